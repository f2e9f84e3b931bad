//! Studs of a two-level grid (docs/fabrication.md, "Joints"): at every A×B node a
//! square stud stands along the surface normal through the gaps of the
//! upper (family A) and the lower (family B) doubled strip; one fastener
//! through each level's two lamellas and the stud holds it. Studs are sawn
//! from bar stock: a cut list, not a sheet part.
//!
//! The stud's section is gap × gap (the profile states no other section, so
//! it can never be larger than the gap). Its middle sits on the surface, so
//! the lamella mid-heights of family A lie `level_offset_mm` (o) above it and
//! those of family B o below.
//!
//! Length rule: the stud passes the full height h of both levels' lamellas,
//! which span o ± h/2 on either side of its middle, so
//!
//! ```text
//! length_mm ≥ 2·o + h
//! ```
//!
//! (the poplar prototype: 2·30 + 60 = 120 mm, exactly its stud).
//!
//! Part frame: x along the stud from its lower end (family B's side, −normal)
//! to its upper end, y across one face, 0 to gap. The fastener holes sit at
//! x = length/2 ∓ o (B, A) on the face's centre line, y = gap/2. The A
//! fastener runs along the A strip's y, the B fastener along the B strip's:
//! at the 90° the studs enforce they are drilled through neighbouring
//! faces, a quarter turn apart about the stud's axis; the 2D part shows
//! both on one face.

use crate::error::{Error, Result};
use crate::fabricate::part::{HoleUse, Part, PartKind};
use crate::profile::{JointSystem, Profile};
use kurbo::Point;

/// Part id of the stud.
pub const STUD_ID: &str = "ST";

/// The studs of a grid: the part and what it takes from bar stock.
#[derive(Debug, Clone, PartialEq)]
pub struct StudCut {
    /// The stud, `count` = number of A×B nodes.
    pub part: Part,
    /// Studs sawn from one bar: n with n·length + (n − 1)·kerf ≤ bar length.
    pub per_bar: u32,
    /// Bars needed for `part.count` studs.
    pub bars: u32,
}

/// How many pieces of `piece_mm` one bar of `bar_mm` yields with a saw
/// kerf of `kerf_mm` between neighbouring pieces: the largest n with
/// n·piece + (n − 1)·kerf ≤ bar (0 when one piece is longer than the bar).
pub fn pieces_per_bar(bar_mm: f64, piece_mm: f64, kerf_mm: f64) -> u32 {
    if piece_mm <= 0.0 || bar_mm < piece_mm {
        return 0;
    }
    // A tiny slack so that an exact fit is not lost to rounding.
    let n = ((bar_mm + kerf_mm) / (piece_mm + kerf_mm) + 1e-9).floor();
    n.min(f64::from(u32::MAX)) as u32
}

/// The studs of a two-level grid with `nodes` A×B nodes: `None` when the
/// joint is not two-level, the profile has no stud, or there are no nodes.
///
/// Errors (one line naming the profile and the part class `ST`): a fastener
/// as wide as the stud or wider (the hole would cut it in two), or as wide
/// as the lamella height; a stud shorter than 2·level offset + lamella
/// height (it would not pass through both levels, see the module doc); a
/// stud longer than the bar it is sawn from.
pub fn studs(profile: &Profile, nodes: usize) -> Result<Option<StudCut>> {
    let Some(stud) = &profile.stud else {
        return Ok(None);
    };
    if profile.joint.system != JointSystem::TwoLevel || nodes == 0 {
        return Ok(None);
    }
    let fail = |what: String| Err(Error::fabrication_part(&profile.source, STUD_ID, what));
    let side = profile.section.gap_mm;
    let h = profile.section.height_mm;
    let o = profile.joint.level_offset_mm;
    let (len, d) = (stud.length_mm, stud.fastener_diameter_mm);
    if d >= side {
        return fail(format!(
            "the {d} mm fastener is as wide as the {side} × {side} mm stud or wider: its hole cuts the stud in two"
        ));
    }
    if d >= h {
        return fail(format!(
            "the {d} mm fastener does not fit the {h} mm lamella height"
        ));
    }
    let need = 2.0 * o + h;
    if len < need - 1e-9 {
        return fail(format!(
            "a {len} mm stud does not pass through both levels: it needs 2 × {o} mm level offset + {h} mm lamella height = {need} mm"
        ));
    }
    // Sawn with the bar group's kerf.
    let kerf_mm = profile.piece_cutting(crate::profile::Piece::Stud).kerf_mm;
    let per_bar = pieces_per_bar(stud.bar_length_mm, len, kerf_mm);
    if per_bar == 0 {
        return fail(format!(
            "a {len} mm stud is longer than the {} mm bar it is sawn from",
            stud.bar_length_mm
        ));
    }
    let count = u32::try_from(nodes).unwrap_or(u32::MAX);
    // By x: family B's level (lower), then family A's.
    let hole = |x: f64| (Point::new(x, 0.5 * side), d, HoleUse::Node);
    let holes = [hole(0.5 * len - o), hole(0.5 * len + o)];
    let part = super::rectangle_part(STUD_ID, PartKind::Stud, count, len, side, &holes);
    Ok(Some(StudCut {
        part,
        per_bar,
        bars: count.div_ceil(per_bar),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabricate::part::FeatureKind;
    use crate::formats::read::profile_file;
    use crate::geom::plane::signed_area_mm2;
    use std::path::Path;

    fn poplar() -> Profile {
        let mut p = profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/poplar-ply-4.yaml"
        )))
        .expect("poplar profile");
        p.source = "poplar.yaml".into();
        p
    }

    #[test]
    fn poplar_studs_are_a_cut_list() {
        let p = poplar();
        let cut = studs(&p, 37).expect("studs").expect("two-level");
        let s = &cut.part;
        assert_eq!((s.id.as_str(), s.kind, s.count), ("ST", PartKind::Stud, 37));
        assert_eq!((s.length_mm, s.height_mm), (120.0, 20.0));
        assert!((signed_area_mm2(&s.outline_part_mm) - 120.0 * 20.0).abs() < 1e-9);
        // Holes at the lamella mid-heights: 60 ∓ 30 mm, on the face's centre line.
        let xs: Vec<f64> = s.features.iter().map(|f| f.center_part_mm.x).collect();
        assert_eq!(xs, [30.0, 90.0]);
        assert!(s.holes_part_mm.is_empty());
        for (f, h) in s.features.iter().zip(&s.hole_polygons()) {
            assert_eq!(f.kind, FeatureKind::Hole);
            assert_eq!(f.hole_use, Some(HoleUse::Node));
            assert_eq!((f.center_part_mm.y, f.width_mm), (10.0, 4.0));
            assert!(signed_area_mm2(h) < 0.0);
            for q in h {
                assert!((q.distance(f.center_part_mm) - 2.0).abs() < 1e-9);
            }
        }
        assert!(s.engraving.is_empty());
        // 2000 mm bars, 0.3 mm kerf: 16 × 120 + 15 × 0.3 = 1924.5 ≤ 2000 < 17 × 120 + 16 × 0.3.
        assert_eq!(cut.per_bar, 16);
        assert_eq!(cut.bars, 3);
    }

    /// A kerf of the bars' own (`stocks.stud.kerf_mm`) is the one the
    /// studs are sawn with: at 10 mm, 16 × 120 + 15 × 10 = 2070 > 2000, so
    /// 15 to a bar (15 × 120 + 14 × 10 = 1940).
    #[test]
    fn studs_are_sawn_with_the_bars_own_kerf() {
        let mut p = poplar();
        let entry = p
            .stocks
            .iter_mut()
            .find(|e| e.piece == crate::profile::Piece::Stud)
            .expect("poplar's stud stock");
        entry.kerf_mm = Some(10.0);
        let cut = studs(&p, 37).expect("studs").expect("two-level");
        assert_eq!((cut.per_bar, cut.bars), (15, 3));
        let cut = studs(&p, 46).expect("studs").expect("two-level");
        assert_eq!((cut.per_bar, cut.bars), (15, 4));
    }

    #[test]
    fn pieces_per_bar_counts_the_kerf_between_pieces() {
        assert_eq!(pieces_per_bar(1000.0, 100.0, 0.0), 10);
        assert_eq!(pieces_per_bar(1000.0, 100.0, 1.0), 9);
        assert_eq!(pieces_per_bar(1009.0, 100.0, 1.0), 10);
        assert_eq!(pieces_per_bar(99.0, 100.0, 1.0), 0);
        assert_eq!(pieces_per_bar(100.0, 100.0, 5.0), 1);
    }

    #[test]
    fn no_studs_without_a_two_level_joint() {
        let steel = profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/steel-1.5.yaml"
        )))
        .expect("steel");
        assert_eq!(studs(&steel, 10).expect("ok"), None);
        assert_eq!(studs(&poplar(), 0).expect("ok"), None);
    }

    #[test]
    fn errors_name_the_stud_class() {
        let msg = |p: &Profile| studs(p, 4).expect_err("must fail").to_string();
        let mut wide = poplar();
        if let Some(s) = wide.stud.as_mut() {
            s.fastener_diameter_mm = 20.0;
        }
        let m = msg(&wide);
        assert!(
            m.starts_with("poplar.yaml: part ST: ") && m.contains("cuts the stud"),
            "{m}"
        );
        let mut short = poplar();
        if let Some(s) = short.stud.as_mut() {
            s.length_mm = 119.0;
        }
        let m = msg(&short);
        assert!(m.contains("both levels") && m.contains("120 mm"), "{m}");
        let mut bar = poplar();
        if let Some(s) = bar.stud.as_mut() {
            s.bar_length_mm = 100.0;
        }
        assert!(msg(&bar).contains("longer than the 100 mm bar"));
        assert!(!msg(&short).contains('\n'));
    }
}
