//! The kit as a strip-packing instance for sparrow (jagua-rs 0.7 JSON):
//! `{name, strip_height, items: [{id, demand, allowed_orientations: [deg…],
//! shape: {type: "simple_polygon", data: [[x, y]…]}}]}`. The strip height is
//! the sheet's width less the margins; every part's outline is grown by
//! half the kerf plus part spacing, so parts that merely touch in sparrow's
//! nest are the right distance apart when cut. Holes are dropped (jagua-rs
//! items have none); slots narrower than the growth close.

use crate::fabricate::Kit;
use crate::nest::outline::grown_outline;
use crate::profile::Profile;
use serde::Serialize;

/// The instance file.
#[derive(Debug, Serialize)]
pub struct Instance {
    /// Instance name (the network's).
    pub name: String,
    /// Usable sheet width, mm.
    pub strip_height: f64,
    /// One per distinct part.
    pub items: Vec<Item>,
}

/// One distinct part.
#[derive(Debug, Serialize)]
pub struct Item {
    /// Index in the kit's parts.
    pub id: usize,
    /// Copies wanted.
    pub demand: u32,
    /// Allowed rotations, degrees.
    pub allowed_orientations: Vec<f64>,
    /// The grown outline.
    pub shape: Shape,
}

/// A polygon shape.
#[derive(Debug, Serialize)]
pub struct Shape {
    /// Always `simple_polygon`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Vertices, counter-clockwise, mm.
    pub data: Vec<[f64; 2]>,
}

/// The instance of a kit for a profile's stock (with several sizes, the
/// strip is as high as the widest size's usable width).
pub fn instance(name: &str, kit: &Kit, profile: &Profile) -> Instance {
    let c = &profile.cutting;
    let d = 0.5 * (c.kerf_mm + c.part_spacing_mm);
    let round = |x: f64| (x * 1e4).round() / 1e4 + 0.0;
    Instance {
        name: name.to_string(),
        strip_height: round(profile.stock.widest_usable_mm(c.edge_margin_mm)),
        items: kit
            .parts
            .iter()
            .enumerate()
            .map(|(i, p)| Item {
                id: i,
                demand: p.count,
                allowed_orientations: c
                    .allowed_rotations_deg
                    .iter()
                    .map(|&r| f64::from(r))
                    .collect(),
                shape: Shape {
                    kind: "simple_polygon".into(),
                    data: grown_outline(p, d)
                        .iter()
                        .map(|q| [round(q.x), round(q.y)])
                        .collect(),
                },
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabricate::part::signed_area_mm2;
    use crate::fabricate::part::{Feature, FeatureKind, Part, PartKind, SlotEdge};
    use kurbo::Point;

    fn part(kind: PartKind, outline: Vec<Point>, features: Vec<Feature>) -> Part {
        Part {
            id: "P".into(),
            kind,
            strip: None,
            lamella: None,
            count: 1,
            length_mm: 100.0,
            height_mm: 50.0,
            station_start_mm: None,
            outline_part_mm: outline,
            holes_part_mm: Vec::new(),
            engraving: Vec::new(),
            features,
        }
    }

    fn rect() -> Vec<Point> {
        vec![
            Point::new(0.0, 0.0),
            Point::new(100.0, 0.0),
            Point::new(100.0, 50.0),
            Point::new(0.0, 50.0),
        ]
    }

    #[test]
    fn a_rectangle_grows_by_d_all_round() {
        let g = grown_outline(&part(PartKind::ShearBlock, rect(), Vec::new()), 2.0);
        assert!((signed_area_mm2(&g) - 104.0 * 54.0).abs() < 1e-9);
        assert!(g.contains(&Point::new(-2.0, -2.0)) && g.contains(&Point::new(102.0, 52.0)));
    }

    #[test]
    fn lamella_notches_narrow_and_close() {
        let slot = |x: f64, w: f64| Feature {
            kind: FeatureKind::Slot,
            hole_use: None,
            node: None,
            crossing: None,
            center_part_mm: Point::new(x, 37.5),
            width_mm: w,
            depth_mm: 25.0,
            edge: Some(SlotEdge::Top),
            angle_range_deg: None,
            station_mm: None,
        };
        let p = part(
            PartKind::Lamella,
            rect(),
            vec![slot(30.0, 10.0), slot(70.0, 3.0)],
        );
        let g = grown_outline(&p, 2.0);
        // The 10 mm slot stays, 6 mm wide, its root 2 mm higher (25 mm below
        // the grown edge); the 3 mm one closes.
        let area = 104.0 * 54.0 - 6.0 * 25.0;
        assert!(
            (signed_area_mm2(&g) - area).abs() < 1e-9,
            "{}",
            signed_area_mm2(&g)
        );
    }
}
