//! Eye plates: the flat plates a bracing cable is pinned to
//! ([`crate::structure::bracing`]), one at each end of every cable, under
//! the bolt of the joint it ends at (the node bolt at an A×B node, the
//! edge bolt at an edge node), on top of the star washer.
//!
//! Geometry (`bracing.eye_plate` of the profile), in the part's frame: an
//! obround `width_mm` (w) wide, its two ends half circles of radius w/2
//! about the two holes' centres, `hole_spacing_mm` (s) apart along x: the
//! bolt's hole (its diameter plus the bolt's hole clearance) at
//! (w/2, w/2), the pin's hole (`pin_hole_mm`) at (w/2 + s, w/2). The
//! outline is `length_mm` = s + w long and w high; its end arcs are
//! polylines whose vertices lie on the arcs and whose chords stray at most
//! [`ARC_TOLERANCE_MM`] inside them (an even number of chords per half
//! circle, so the tips at x = 0 and x = s + w are vertices and the
//! bounding box is exact). The plate turns about its bolt to point along
//! its cable, so one part serves every cable end on bolts of one diameter:
//! `EP8` for an M8 bolt, its count the cable ends there.
//!
//! Several cables ending at one joint stack their plates under its bolt:
//! the bolt's grip grows by a plate thickness for each
//! ([`super::hardware`]).

use super::part::{Feature, FeatureKind, HoleUse, Part, PartKind, ARC_TOLERANCE_MM};
use crate::profile::EyePlate;
use kurbo::Point;

/// The part id of the eye plates on bolts of `bolt_diameter_mm`: `EP8`,
/// `EP10`.
pub fn eye_plate_id(bolt_diameter_mm: f64) -> String {
    format!("EP{}", crate::profile::groups::trim_mm(bolt_diameter_mm))
}

/// Chords of a half circle of `radius_mm` whose chords stray at most
/// `tolerance_mm` inside it: even, at least 4.
fn half_circle_chords(radius_mm: f64, tolerance_mm: f64) -> usize {
    let half_angle = (1.0 - (tolerance_mm / radius_mm).min(1.0)).acos();
    let n = (std::f64::consts::FRAC_PI_2 / half_angle.max(1e-6)).ceil() as usize;
    (2 * n).clamp(4, 720)
}

/// The obround's outline, counter-clockwise from the bottom edge's start,
/// in the part frame (see the module doc).
pub fn eye_plate_outline(plate: &EyePlate) -> Vec<Point> {
    let r = 0.5 * plate.width_mm;
    let (bolt, pin) = (Point::new(r, r), Point::new(r + plate.hole_spacing_mm, r));
    let n = half_circle_chords(r, ARC_TOLERANCE_MM);
    let arc = |c: Point, from: f64| {
        (0..=n).map(move |k| {
            let a = from + std::f64::consts::PI * k as f64 / n as f64;
            Point::new(c.x + r * a.cos(), c.y + r * a.sin())
        })
    };
    let half_pi = std::f64::consts::FRAC_PI_2;
    arc(pin, -half_pi).chain(arc(bolt, half_pi)).collect()
}

/// The eye plate for bolts of `bolt_diameter_mm` with holes
/// `hole_clearance_mm` wider, `count` times.
pub fn eye_plate_part(
    plate: &EyePlate,
    bolt_diameter_mm: f64,
    hole_clearance_mm: f64,
    count: u32,
) -> Part {
    let r = 0.5 * plate.width_mm;
    let hole = |x: f64, d: f64, u: HoleUse| Feature {
        kind: FeatureKind::Hole,
        hole_use: Some(u),
        node: None,
        crossing: None,
        center_part_mm: Point::new(x, r),
        width_mm: d,
        depth_mm: 0.0,
        edge: None,
        angle_range_deg: None,
        station_mm: None,
    };
    Part {
        id: eye_plate_id(bolt_diameter_mm),
        kind: PartKind::EyePlate,
        strip: None,
        lamella: None,
        count,
        length_mm: plate.hole_spacing_mm + plate.width_mm,
        height_mm: plate.width_mm,
        station_start_mm: None,
        outline_part_mm: eye_plate_outline(plate),
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features: vec![
            hole(r, bolt_diameter_mm + hole_clearance_mm, HoleUse::Node),
            hole(
                r + plate.hole_spacing_mm,
                plate.pin_hole_mm,
                HoleUse::CablePin,
            ),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::plane::signed_area_mm2;

    fn plate() -> EyePlate {
        EyePlate {
            thickness_mm: 4.0,
            width_mm: 24.0,
            hole_spacing_mm: 30.0,
            pin_hole_mm: 6.5,
            yield_mpa: None,
        }
    }

    /// The outline is the obround: every vertex on its end circles (the
    /// straight sides join them), counter-clockwise, its bounding box
    /// s + w by w from the origin, its area within the chords' loss of
    /// w·s + π·(w/2)² (each chord of a half circle loses less than
    /// tolerance × its length).
    #[test]
    fn outline_is_the_obround() {
        let p = plate();
        let out = eye_plate_outline(&p);
        let r = 12.0;
        for q in &out {
            // On the end circle of its side: the bolt's up to x = w/2,
            // the pin's from x = w/2 + s (the straight sides are chords).
            let centre = if q.x <= r + 1e-9 {
                Point::new(r, r)
            } else {
                Point::new(r + 30.0, r)
            };
            assert!((q.distance(centre) - r).abs() < 1e-9, "{q:?}");
            assert!(q.x <= r + 1e-9 || q.x >= r + 30.0 - 1e-9, "{q:?}");
        }
        let xs = out.iter().map(|q| q.x);
        assert!((xs.clone().fold(f64::INFINITY, f64::min)).abs() < 1e-9);
        assert!((xs.fold(f64::NEG_INFINITY, f64::max) - 54.0).abs() < 1e-9);
        let area = signed_area_mm2(&out);
        let exact = 24.0 * 30.0 + std::f64::consts::PI * r * r;
        assert!(area > 0.0, "counter-clockwise");
        assert!(area < exact && exact - area < ARC_TOLERANCE_MM * 2.0 * std::f64::consts::PI * r);
    }

    /// The part: id by bolt, holes at the two centres, bolt hole with its
    /// clearance, the pin's hole marked as such.
    #[test]
    fn part_holes_and_id() {
        let part = eye_plate_part(&plate(), 8.0, 1.0, 6);
        assert_eq!((part.id.as_str(), part.count), ("EP8", 6));
        assert_eq!((part.length_mm, part.height_mm), (54.0, 24.0));
        let holes: Vec<(f64, f64, f64)> = part
            .round_holes()
            .into_iter()
            .map(|(c, r)| (c.x, c.y, 2.0 * r))
            .collect();
        assert_eq!(holes, vec![(12.0, 12.0, 9.0), (42.0, 12.0, 6.5)]);
        assert_eq!(part.features[1].hole_use, Some(HoleUse::CablePin));
        assert_eq!(eye_plate_id(10.0), "EP10");
    }

    /// EN 1993-1-8 Table 3.9 by hand ([`EyePlate::pin_resistance_n`]): 4 mm S355 plate 24 mm wide, 6.5 mm
    /// pin hole: a = (24 − 6.5)/2 = 8.75, a − 2·6.5/3 = 4.4167, F_Rd =
    /// 2·4·355·4.4167 = 12 543 N. A 3 mm rim beside a 12 mm hole leaves
    /// nothing: 0.
    #[test]
    fn pin_resistance_by_hand() {
        let f = plate().pin_resistance_n(355.0, 1.0);
        assert!((f - 2.0 * 4.0 * 355.0 * (8.75 - 13.0 / 3.0)).abs() < 1e-9);
        assert!((f - 12_543.33).abs() < 0.01, "{f}");
        let thin = EyePlate {
            width_mm: 18.0,
            pin_hole_mm: 12.0,
            ..plate()
        };
        assert_eq!(thin.pin_resistance_n(355.0, 1.0), 0.0);
    }
}
