//! Stock from the profile: several sheet sizes with prices and
//! count limits, and coil cut to length. Figures are held to values
//! computed by hand or by brute force over sheet mixes, not read back from
//! the nest.

use crate::support::{self, root};
use kurbo::Point;
use lamella::fabricate::part::{Part, PartKind};
use lamella::fabricate::{fabricate, Kit, KitSummary};
use lamella::formats::read::profile_file;
use lamella::formats::read::{read_network, ReadOptions};
use lamella::nest::{check_nest, nest, Nest};
use lamella::profile::Profile;
use lamella::{analyze, AnalysisOptions};
use std::path::Path;

/// The steel profile's text with its `stock:` section replaced.
fn steel_with(stock: &str) -> String {
    let s = std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).unwrap();
    let a = s.find("stock:\n").unwrap();
    let b = s.find("cutting:\n").unwrap();
    format!("{}{stock}{}", &s[..a], &s[b..])
}

fn parse(text: &str) -> lamella::Result<Profile> {
    profile_file::parse(text, Path::new("test.yaml"))
}

/// Large 3000 × 1500 (27 lanes of 2983.2 mm for 50 mm lamellas 3.2 mm
/// apart) and small 2000 × 1000 (18 lanes of 1983.2 mm), with prices and
/// limits.
fn two_sizes(large: f64, small: f64, limits: (Option<u32>, Option<u32>)) -> Profile {
    let limit = |n: Option<u32>| n.map(|n| format!(", max_count: {n}")).unwrap_or_default();
    parse(&steel_with(&format!(
        "stock:\n  kind: sheet\n  currency: EUR\n  sizes:\n    \
         - {{length_mm: 3000, width_mm: 1500, price_per_unit: {large}{}}}\n    \
         - {{length_mm: 2000, width_mm: 1000, price_per_unit: {small}{}}}\n",
        limit(limits.0),
        limit(limits.1)
    )))
    .unwrap()
}

/// A kit of lamella rectangles: (length, count) each, 50 mm high.
fn lamellas(parts: &[(f64, u32)]) -> Kit {
    let parts = parts
        .iter()
        .enumerate()
        .map(|(k, &(len, count))| Part {
            id: format!("L{k}"),
            kind: PartKind::Lamella,
            strip: None,
            lamella: Some(1),
            count,
            length_mm: len,
            height_mm: 50.0,
            station_start_mm: Some(0.0),
            outline_part_mm: vec![
                Point::new(0.0, 0.0),
                Point::new(len, 0.0),
                Point::new(len, 50.0),
                Point::new(0.0, 50.0),
            ],
            holes_part_mm: Vec::new(),
            engraving: Vec::new(),
            features: Vec::new(),
        })
        .collect();
    Kit {
        parts,
        summary: KitSummary::default(),
        warnings: Vec::new(),
    }
}

fn sheets_of(n: &Nest, stock: &str) -> usize {
    n.sheets.iter().filter(|s| s.stock == stock).count()
}

#[test]
fn every_stock_form_reads_and_writes_back() {
    for stock in [
        "stock:\n  kind: sheet\n  length_mm: 3000\n  width_mm: 1500\n  max_count: 4\n",
        "stock:\n  kind: sheet\n  sizes:\n    - {name: large, length_mm: 3000, width_mm: 1500, max_count: 2}\n    - {length_mm: 2000, width_mm: 1000}\n",
        "stock:\n  kind: coil\n  width_mm: 130\n  price_per_m: 12.5\n  currency: EUR\n  length_step_mm: 10\n",
        "stock:\n  kind: coil\n  width_mm: 130\n  length_mm: 6000\n  price_per_unit: 40\n",
    ] {
        let text = steel_with(stock);
        let file: profile_file::ProfileFile = serde_yaml::from_str(&text).unwrap();
        let p = parse(&text).unwrap_or_else(|e| panic!("{stock}: {e}"));
        assert_eq!(profile_file::ProfileFile::from(&p), file, "{stock}");
    }
    let p = two_sizes(95.0, 45.0, (None, Some(3)));
    assert_eq!(p.stock.sizes.len(), 2);
    assert_eq!(p.stock.sizes[1].label(), "2000 × 1000");
    assert_eq!(p.stock.sizes[1].max_count, Some(3));
    // The longest usable length is what a lamella may be.
    assert_eq!(p.stock.longest_usable_mm(10.0, 50.0), 2980.0);
    let mixed = support::profile("steel-1.5-mixed");
    assert_eq!(mixed.stock.sizes.len(), 2);
    assert!(mixed.stock.priced());
}

#[test]
fn bad_stock_fields_are_named_in_one_line() {
    let size = |extra: &str| {
        format!(
            "stock:\n  kind: sheet\n  sizes:\n    - {{length_mm: 3000, width_mm: 1500, price_per_unit: 95}}\n    - {{length_mm: 2000, width_mm: 1000{extra}}}\n"
        )
    };
    let cases: Vec<(String, &[&str])> = vec![
        (size(""), &["stock.sizes[1].price_per_unit", "every size or for none"]),
        (size(", price_per_unit: 45, max_count: 0"), &["stock.sizes[1].max_count", "at least 1"]),
        (size(", price_per_unit: -45"), &["stock.sizes[1].price_per_unit", "zero or more"]),
        (size(", price_per_unit: 45, colour: red"), &["unknown field `colour`"]),
        (
            "stock:\n  kind: sheet\n  sizes:\n    - {length_mm: 3000, width_mm: -1}\n".into(),
            &["stock.sizes[0].width_mm", "positive"],
        ),
        (
            "stock:\n  kind: sheet\n  sizes:\n    - {length_mm: 3000, width_mm: 1500}\n    - {length_mm: 3000, width_mm: 1500}\n".into(),
            &["stock.sizes[1].length_mm", "stock.sizes[0] again"],
        ),
        (
            "stock:\n  kind: sheet\n  sizes:\n    - {length_mm: 3000, width_mm: 40}\n".into(),
            &["stock.sizes[0].width_mm", "narrower than a lamella"],
        ),
        (
            "stock:\n  kind: sheet\n  length_mm: 3000\n  sizes:\n    - {length_mm: 3000, width_mm: 1500}\n".into(),
            &["stock.length_mm", "per size"],
        ),
        ("stock:\n  kind: sheet\n  sizes: []\n".into(), &["stock.sizes", "at least one"]),
        ("stock:\n  kind: sheet\n  width_mm: 1500\n".into(), &["stock.length_mm", "missing"]),
        (
            "stock:\n  kind: sheet\n  length_mm: 3000\n  width_mm: 1500\n  price_per_m: 3\n".into(),
            &["stock.price_per_m", "coil"],
        ),
        (
            "stock:\n  kind: coil\n  sizes:\n    - {length_mm: 3000, width_mm: 1500}\n".into(),
            &["stock.sizes", "one width"],
        ),
        ("stock:\n  kind: coil\n  length_mm: 3000\n".into(), &["stock.width_mm", "missing"]),
        (
            "stock:\n  kind: coil\n  width_mm: 130\n  price_per_unit: 40\n".into(),
            &["stock.price_per_unit", "per piece"],
        ),
        (
            "stock:\n  kind: coil\n  width_mm: 130\n  max_count: 3\n".into(),
            &["stock.max_count", "pieces"],
        ),
        (
            "stock:\n  kind: coil\n  width_mm: 130\n  length_mm: 6000\n  price_per_unit: 40\n  price_per_m: 7\n".into(),
            &["stock.price_per_m", "not both"],
        ),
        (
            "stock:\n  kind: coil\n  width_mm: 130\n  length_step_mm: 0\n".into(),
            &["stock.length_step_mm", "positive"],
        ),
    ];
    for (stock, fragments) in cases {
        let e = parse(&steel_with(&stock)).unwrap_err().to_string();
        assert!(!e.contains('\n'), "{e}");
        for f in fragments {
            assert!(e.contains(f), "{stock}: `{f}` not in {e}");
        }
    }
}

/// Lamellas of 900 mm (903.2 mm with the gap): 3 to a large lane, 81 to a
/// large sheet; 2 to a small lane, 36 to a small sheet. The cheapest mix
/// for n lamellas, by brute force over the number of large sheets.
fn cheapest(n: u32, large: f64, small: f64, limits: (u32, u32)) -> Option<f64> {
    (0..=limits.0.min(n.div_ceil(81)))
        .filter_map(|l| {
            let s = n.saturating_sub(81 * l).div_ceil(36);
            (s <= limits.1).then(|| f64::from(l) * large + f64::from(s) * small)
        })
        .min_by(f64::total_cmp)
}

#[test]
fn small_sheets_win_where_they_hold_the_kit_for_less() {
    // Large is the better value per area (85 / 4.41 m² < 40 / 1.94 m²),
    // but 144 lamellas fill exactly 4 small sheets (160) and need 2 large
    // ones (170) or 1 large and 2 small (165).
    let p = two_sizes(85.0, 40.0, (None, None));
    let kit = lamellas(&[(900.0, 144)]);
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    assert_eq!(cheapest(144, 85.0, 40.0, (99, 99)), Some(160.0));
    assert_eq!(n.summary.cost, Some(160.0));
    assert_eq!(sheets_of(&n, "2000 × 1000"), 4);
    assert_eq!(n.summary.sheets_used, 4);
    assert!(n.summary.cost_bound.unwrap() <= 160.0);
    // Every size stated per sheet, with its price.
    assert!(n.sheets.iter().all(|s| s.price_per_unit == Some(40.0)));
    assert_eq!(n.stock_used.len(), 1);
    assert_eq!(n.stock_used[0].cost, Some(160.0));
    // 84 lamellas at 70 for a large sheet: one large and one small (110)
    // beat three small (120) and two large (140).
    let p = two_sizes(70.0, 40.0, (None, None));
    let kit = lamellas(&[(900.0, 84)]);
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    assert_eq!(n.summary.cost, Some(110.0));
    assert_eq!(
        (sheets_of(&n, "3000 × 1500"), sheets_of(&n, "2000 × 1000")),
        (1, 1)
    );
}

/// For every kit of 1 to 300 such lamellas and three price ratios, the
/// nest's cost is the brute-force optimum.
#[test]
fn uniform_kits_cost_the_brute_force_optimum() {
    let mut worse = Vec::new();
    for (large, small) in [(95.0, 45.0), (85.0, 40.0), (70.0, 40.0)] {
        let p = two_sizes(large, small, (None, None));
        for count in 1..=300 {
            let kit = lamellas(&[(900.0, count)]);
            let n = nest(&kit, &p).unwrap();
            assert_eq!(check_nest(&kit, &n, &p), Ok(()));
            let best = cheapest(count, large, small, (999, 999)).unwrap();
            let cost = n.summary.cost.unwrap();
            assert!(
                cost >= best - 1e-9,
                "{count}: {cost} below the optimum {best}"
            );
            if cost > best + 1e-9 {
                worse.push(format!("{count} at {large}/{small}: {cost} vs {best}"));
            }
        }
    }
    assert!(worse.is_empty(), "{worse:?}");
}

#[test]
fn a_count_limit_brings_in_the_second_size() {
    // Small is the better buy here (4 × 40 = 160), but only 2 are in stock:
    // 1 large + 2 small (165) beat 2 large (170).
    let p = two_sizes(85.0, 40.0, (None, Some(2)));
    let kit = lamellas(&[(900.0, 144)]);
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    assert_eq!(cheapest(144, 85.0, 40.0, (99, 2)), Some(165.0));
    assert_eq!(n.summary.cost, Some(165.0));
    assert_eq!(sheets_of(&n, "2000 × 1000"), 2);
    assert_eq!(sheets_of(&n, "3000 × 1500"), 1);
    // Sheets in size order: the large first.
    assert_eq!(n.sheets[0].stock, "3000 × 1500");
    assert_eq!(n.sheets[0].id, "S01");
}

#[test]
fn count_limits_too_small_are_a_one_line_error_saying_what_is_missing() {
    // 1 large (81) + 1 small (36) hold 117 of 144: 27 lamellas, 24.3 m, left.
    let p = two_sizes(85.0, 40.0, (Some(1), Some(1)));
    let kit = lamellas(&[(900.0, 144)]);
    let e = nest(&kit, &p).unwrap_err().to_string();
    assert!(!e.contains('\n'), "{e}");
    for f in [
        "stock",
        "max_count 1 of 3000 × 1500, 1 of 2000 × 1000",
        "27 lamella(s), 24.3 m",
        "1 more sheet(s) of",
    ] {
        assert!(e.contains(f), "`{f}` not in {e}");
    }
    // The single-size form's limit too.
    let p = parse(&steel_with(
        "stock:\n  kind: sheet\n  length_mm: 3000\n  width_mm: 1500\n  max_count: 1\n",
    ))
    .unwrap();
    let e = nest(&kit, &p).unwrap_err().to_string();
    assert!(e.contains("63 lamella(s), 56.7 m"), "{e}");
}

#[test]
fn a_lamella_longer_than_the_small_size_goes_on_the_large_one() {
    // 2500 mm fits only the large lanes; the 900 mm ones fill the rest.
    let p = two_sizes(85.0, 40.0, (None, None));
    let kit = lamellas(&[(2500.0, 3), (900.0, 10)]);
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    // 3 lanes of 2500 + 4 lanes of 900 × 3 (the last 1): one large sheet,
    // 85; no mix is cheaper (the long ones need a large sheet).
    assert_eq!(n.summary.cost, Some(85.0));
    assert_eq!(n.summary.sheets_used, 1);
    // Longer than every size: the existing error naming the part.
    let kit = lamellas(&[(2990.0, 1)]);
    let e = nest(&kit, &p).unwrap_err().to_string();
    assert!(e.contains("part L0") && e.contains("does not fit"), "{e}");
}

/// Coil 130 mm wide: 110 mm usable, 2 lanes of 50 mm lamellas. Lamellas of
/// 1500, 1500, 1000, 1000, 1000 mm with the gap (1496.8 and 996.8 mm):
/// the longest-first greedy gives lanes of 3500 and 2500; the best split
/// is 1500 + 1500 | 1000 + 1000 + 1000, 3000 each: a lane of
/// 3000 − 3.2 = 2996.8 mm of cut, plus the margins 2 × 10 = 3016.8 mm,
/// 3020 mm in 10 mm steps; at 12.50 EUR/m, 37.75 EUR.
#[test]
fn coil_is_cut_to_the_hand_computed_lane_length() {
    let p = parse(&steel_with(
        "stock:\n  kind: coil\n  width_mm: 130\n  price_per_m: 12.5\n  currency: EUR\n  length_step_mm: 10\n",
    ))
    .unwrap();
    let kit = lamellas(&[(1496.8, 2), (996.8, 3)]);
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    let s = &n.summary;
    assert_eq!(s.sheets_used, 1);
    assert_eq!(s.lanes_per_sheet, 2);
    assert_eq!(s.lanes_used, 2);
    assert_eq!(s.length_used_mm, Some(3020.0));
    assert_eq!(n.sheets[0].length_mm, 3020.0);
    assert_eq!(n.sheets[0].width_mm, 130.0);
    assert!((s.length_bound_mm.unwrap() - 3016.8).abs() < 1e-6);
    assert!((s.cost.unwrap() - 37.75).abs() < 1e-9);
    assert_eq!(n.sheets[0].stock, "coil 130");
    // With 2000 mm pieces (lanes of 1983.2): five lanes, three pieces, each
    // cut to its longest lane: 1516.8 → 1520, 1016.8 → 1020 twice.
    let p = parse(&steel_with(
        "stock:\n  kind: coil\n  width_mm: 130\n  length_mm: 2000\n  price_per_m: 12.5\n  length_step_mm: 10\n",
    ))
    .unwrap();
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    assert_eq!(n.summary.sheets_used, 3);
    assert_eq!(n.summary.length_used_mm, Some(3560.0));
    let lengths: Vec<f64> = n.sheets.iter().map(|s| s.length_mm).collect();
    assert_eq!(lengths, [1520.0, 1020.0, 1020.0]);
    // A coil never splices: the lamellas of a 4 m network stay whole.
    let net = read_network(
        &root().join("samples/enneper-4m.yaml"),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let coil = parse(&steel_with(
        "stock:\n  kind: coil\n  width_mm: 1500\n  price_per_m: 60\n",
    ))
    .unwrap();
    let kit = fabricate(&net, &an, &coil, None, Default::default()).unwrap();
    assert!(kit.parts.iter().all(|p| p.kind != PartKind::SplicePlate));
    let n = nest(&kit, &coil).unwrap();
    assert_eq!(check_nest(&kit, &n, &coil), Ok(()));
    let s = &n.summary;
    assert!(s.length_used_mm.unwrap() >= s.length_bound_mm.unwrap());
    assert!(s.cost.unwrap() >= s.cost_bound.unwrap());
}

/// Every buildable sample with the mixed-size steel profile: the
/// invariants, at most the single size's cost, splices at the longest
/// size, deterministic.
#[test]
fn shipped_samples_nest_on_two_sizes_within_the_rules() {
    let mixed = support::profile("steel-1.5-mixed");
    let single = support::profile("steel-1.5");
    let small = parse(&steel_with(
        "stock:\n  kind: sheet\n  length_mm: 2000\n  width_mm: 1000\n  price_per_unit: 45\n",
    ))
    .unwrap();
    for sample in support::BUILDABLE_SAMPLES {
        let (net, an) = support::analysed_sample(sample);
        let kit = fabricate(&net, &an, &mixed, None, Default::default()).unwrap();
        // The same parts as with the large size alone (splices at 2980 mm).
        let kit_single = fabricate(&net, &an, &single, None, Default::default()).unwrap();
        assert_eq!(kit.parts, kit_single.parts, "{sample}");
        let n = nest(&kit, &mixed).unwrap();
        assert_eq!(check_nest(&kit, &n, &mixed), Ok(()), "{sample}");
        let s = &n.summary;
        assert!(s.sheets_used >= s.lower_bound_sheets, "{sample}");
        assert!(s.cost.unwrap() >= s.cost_bound.unwrap(), "{sample}");
        let alone = nest(&kit, &single).unwrap().summary.cost.unwrap();
        assert!(s.cost.unwrap() <= alone, "{sample}: {:?} > {alone}", s.cost);
        let total: f64 = n.sheets.iter().map(|s| s.price_per_unit.unwrap()).sum();
        assert!((total - s.cost.unwrap()).abs() < 1e-9);
        assert_eq!(
            nest(&kit, &mixed).unwrap().sheets,
            n.sheets,
            "{sample}: deterministic"
        );
        // With only the small size, more lamella pieces (splices at 1980).
        if let Ok(k) = fabricate(&net, &an, &small, None, Default::default()) {
            let pieces = |k: &Kit| {
                k.parts
                    .iter()
                    .filter(|p| p.kind == PartKind::Lamella)
                    .count()
            };
            assert!(pieces(&k) >= pieces(&kit), "{sample}");
        }
    }
}
